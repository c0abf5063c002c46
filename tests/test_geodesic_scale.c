/* test_geodesic_scale.c - geodesic results do not depend on the unit or the position of the
 * coordinates (once a square at 1e80 gave a `proven` path 41% long, spot at 1e60
 * asymmetric `proven` paths, fields 3.5% off from 1e55 up and 1e-60 down, all zeros at 1e-300).
 * The corpus's spot and a closed holed plate, scaled by 10^e for e in -150..150 and by 2^k, and
 * translated about a thousand diameters from the origin: fields (from a vertex and from a face
 * point), distances at surface points and paths by every method (with and without the exact
 * check) must equal the unscaled ones divided by the scale to 1e-12, keep their status and
 * label, and no path is `proven` unless its length is the field's distance. (Paths of the
 * straightener and the relaxation on the plate, where equally long edge paths abound, may end in
 * another geodesic: see compare.) Beyond +-1e150 the
 * solver is refused (TG_ERR_UNSUPPORTED), never answers. Then sampling, Voronoi cells, isolines,
 * routes through waypoints and distance matrices on spot scaled by 2^+-330, 2^+-490 and 1e+-100
 * (test_more_commands). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tg_test.h"
#include "tg_test_path.h"
#include "tg_test_plate.h"

#define PAIRS 6
#define RELAX_PAIR 4 /* a pair of face points, the relaxation's quickest of the six */
#define REL 1e-12
/* A proven path is the exact path: its length is the field's distance within the path module's
 * margin for "proven" (1e-9 relative). */
#define PROVEN_REL 1e-9

typedef struct answers {
    double* field_v;   /* field from a vertex, at every vertex */
    double* field_f;   /* field from a face point, at every vertex */
    double at[PAIRS];  /* field_at from[i] -> to[i] */
    double len[PAIRS][4][2];      /* path length per method, certify off / on */
    int status[PAIRS][4][2];
    int global[PAIRS][4][2];
} answers;

typedef struct scene {
    const char* name;
    tg_mesh* unit;       /* coordinates rounded to multiples of 2^-32 of `size` (see quantized) */
    double size;         /* the power of two above the largest coordinate's magnitude */
    double extent;       /* the largest coordinate's magnitude */
    tg_surface_point src_v, src_f;
    tg_surface_point from[PAIRS], to[PAIRS];
    answers ref;
    bool tied;           /* edge paths of equal length abound (see compare) */
    int variants, worst_e, other_geodesic;
    double worst;        /* the largest relative difference seen */
} scene;

/* The mesh with its coordinates rounded to multiples of 2^-32 of its size: any translation by a
 * multiple of 2^10 sizes is then exact, so the translated mesh differs from the unit one only by
 * the rounding of the final scaling. */
static tg_mesh* quantized(const tg_mesh* m, double* out_size, double* out_extent)
{
    const tg_mesh_report* r = tg_mesh_get_report(m);
    double ext = 0.0;
    for (int k = 0; k < 3; ++k) ext = fmax(ext, fmax(fabs(r->bbox_min[k]), fabs(r->bbox_max[k])));
    int e;
    frexp(ext, &e);
    double size = ldexp(1.0, e), q = ldexp(size, -32);
    size_t nv = tg_mesh_vertex_count(m);
    double* xyz = malloc(3 * nv * sizeof *xyz);
    const double* p = tg_mesh_positions(m);
    for (size_t i = 0; i < 3 * nv; ++i) xyz[i] = nearbyint(p[i] / q) * q;
    tg_mesh* out = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tg_mesh_triangles(m), tg_mesh_face_count(m), NULL, NULL, &out), TG_OK);
    free(xyz);
    *out_size = size;
    *out_extent = ext;
    return out;
}

/* The mesh x -> s (x + t) (same faces); x + t is exact (see quantized). */
static tg_mesh* transformed(const tg_mesh* m, double s, double t)
{
    size_t nv = tg_mesh_vertex_count(m);
    double* xyz = malloc(3 * nv * sizeof *xyz);
    const double* p = tg_mesh_positions(m);
    static const double dir[3] = {1.0, -2.0, 4.0};
    for (size_t i = 0; i < 3 * nv; ++i) xyz[i] = s * (p[i] + dir[i % 3] * t);
    tg_mesh* out = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tg_mesh_triangles(m), tg_mesh_face_count(m), NULL, NULL, &out), TG_OK);
    free(xyz);
    return out;
}

/* Every answer of the scene's queries on mesh m (NULL answers: only the solver's refusal is
 * checked by the caller). Each proven path is checked against the field's distance here. */
static tg_status compute(const scene* sc, const tg_mesh* m, answers* a)
{
    tg_geodesic* g = NULL;
    tg_status st = tg_geodesic_create(m, NULL, &g);
    if (st != TG_OK) return st;
    tg_geodesic_workspace* ws = NULL;
    tg_path* path = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &path), TG_OK);
    CHECK_STATUS(tg_geodesic_field(g, ws, &sc->src_v, 1, NULL, a->field_v, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_field(g, ws, &sc->src_f, 1, NULL, a->field_f, NULL), TG_OK);
    for (int i = 0; i < PAIRS; ++i) {
        CHECK_STATUS(tg_geodesic_field_at(g, ws, &sc->from[i], 1, &sc->to[i], 1, NULL, &a->at[i], NULL, NULL), TG_OK);
        for (int k = 0; k < 4; ++k) {
            for (int c = 0; c < 2; ++c) {
                if (tg_test_path_methods[k] == TG_PATH_RELAX && i != RELAX_PAIR) { /* 100x slower: one pair */
                    a->len[i][k][c] = 0.0, a->status[i][k][c] = a->global[i][k][c] = 0;
                    continue;
                }
                if (k == 0 && c == 1) { /* exact: certify changes nothing */
                    a->len[i][k][c] = a->len[i][k][0], a->status[i][k][c] = a->status[i][k][0];
                    a->global[i][k][c] = a->global[i][k][0];
                    continue;
                }
                tg_path_options o;
                memset(&o, 0, sizeof o);
                o.method = tg_test_path_methods[k];
                o.certify = c ? TG_PATH_CERTIFY_ON : TG_PATH_CERTIFY_OFF;
                CHECK_STATUS(tg_geodesic_path(g, ws, &sc->from[i], &sc->to[i], &o, path), TG_OK);
                tg_path_view v;
                tg_path_get_view(path, &v);
                a->len[i][k][c] = v.length, a->status[i][k][c] = (int)v.status, a->global[i][k][c] = (int)v.global;
                CHECK_MSG(v.global != TG_PATH_PROVEN || fabs(v.length - a->at[i]) <= PROVEN_REL * a->at[i],
                          "%s pair %d %s certify %d: proven at %.17g, the field says %.17g", sc->name, i,
                          tg_test_method_name(tg_test_path_methods[k]), c, v.length, a->at[i]);
            }
        }
    }
    tg_path_destroy(path);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    return TG_OK;
}

/* got (on the mesh scaled by s) against want (unit mesh): |got / s - want| <= REL want + slack,
 * slack the bound of what the rounding of the input coordinates can change (0 when scaled only). */
static bool agrees(scene* sc, double got, double want, double s, double slack, int e)
{
    double u = got / s;
    if (isinf(want)) return isinf(got);
    double diff = fabs(u - want);
    if (want > 0.0 && diff / want > sc->worst && diff > slack) sc->worst = diff / want, sc->worst_e = e;
    return diff <= REL * want + slack;
}

static void compare(scene* sc, const answers* a, size_t nv, double s, double slack, int e, const char* how)
{
    const answers* r = &sc->ref;
    int bad_v = 0, bad_f = 0;
    size_t first = 0;
    for (size_t v = 0; v < nv; ++v) {
        if (!agrees(sc, a->field_v[v], r->field_v[v], s, slack, e) && bad_v++ == 0) first = v;
        if (!agrees(sc, a->field_f[v], r->field_f[v], s, slack, e)) bad_f++;
    }
    CHECK_MSG(bad_v == 0 && bad_f == 0, "%s %s: %d + %d field values off (vertex %zu: %.17g vs %.17g)", sc->name, how,
              bad_v, bad_f, first, a->field_v[first] / s, r->field_v[first]);
    for (int i = 0; i < PAIRS; ++i) {
        CHECK_MSG(agrees(sc, a->at[i], r->at[i], s, slack, e), "%s %s pair %d: field_at %.17g vs %.17g", sc->name, how,
                  i, a->at[i] / s, r->at[i]);
        for (int k = 0; k < 4; ++k)
            for (int c = 0; c < 2; ++c) {
                /* On the plate many edge paths are exactly as long (a grid); which one A* keeps,
                 * and so which geodesic the straightener or the relaxation ends in, turns on the
                 * last bit of the input. Such a path must still be no shorter than the exact
                 * distance and keep its status and label; it is counted, not failed. */
                bool local = !c && (tg_test_path_methods[k] == TG_PATH_STRAIGHTEN ||
                                    tg_test_path_methods[k] == TG_PATH_RELAX);
                double worst = sc->worst;
                int worst_e = sc->worst_e;
                if (sc->tied && local && !agrees(sc, a->len[i][k][c], r->len[i][k][c], s, slack, e) &&
                    a->len[i][k][c] / s >= r->at[i] * (1.0 - REL) && a->status[i][k][c] == r->status[i][k][c] &&
                    a->global[i][k][c] == r->global[i][k][c]) {
                    sc->other_geodesic++;
                    sc->worst = worst, sc->worst_e = worst_e; /* not a difference of the same path */
                    continue;
                }
                CHECK_MSG(agrees(sc, a->len[i][k][c], r->len[i][k][c], s, slack, e) &&
                              a->status[i][k][c] == r->status[i][k][c] && a->global[i][k][c] == r->global[i][k][c],
                          "%s %s pair %d %s certify %d: length %.17g (%s, %s) vs %.17g (%s, %s)", sc->name, how, i,
                          tg_test_method_name(tg_test_path_methods[k]), c, a->len[i][k][c] / s,
                          tg_path_status_name((tg_path_status)a->status[i][k][c]),
                          a->global[i][k][c] == TG_PATH_PROVEN ? "proven" : "unproven", r->len[i][k][c],
                          tg_path_status_name((tg_path_status)r->status[i][k][c]),
                          r->global[i][k][c] == TG_PATH_PROVEN ? "proven" : "unproven");
            }
    }
}

static void alloc_answers(answers* a, size_t nv)
{
    a->field_v = malloc(nv * sizeof(double));
    a->field_f = malloc(nv * sizeof(double));
}

static void pick_points(scene* sc, uint64_t seed)
{
    size_t nv = tg_mesh_vertex_count(sc->unit), nf = tg_mesh_face_count(sc->unit);
    tg_rng r = {seed};
    sc->src_v = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
    sc->src_f = random_face_point(&r, nf);
    for (int i = 0; i < PAIRS; ++i) {
        /* half vertex pairs (ties between paths are most likely there), half face points */
        if (i % 2 == 0) {
            sc->from[i] = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
            sc->to[i] = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
        } else {
            sc->from[i] = random_face_point(&r, nf);
            sc->to[i] = random_face_point(&r, nf);
        }
    }
}

static void run_scene(scene* sc)
{
    size_t nv = tg_mesh_vertex_count(sc->unit);
    alloc_answers(&sc->ref, nv);
    CHECK_STATUS(compute(sc, sc->unit, &sc->ref), TG_OK);
    answers a;
    alloc_answers(&a, nv);
    /* the full suite every 10th exponent (50th under the sanitizers); the fast one every 50th
     * (75th): both ends of the range (+-150) and the unit mesh (0) always */
    const int step = TG_TEST_DEPTH(TG_TEST_WORK(10, 50), TG_TEST_WORK(50, 75));
    for (int e = -150; e <= 150; e += step) {
        double s = pow(10.0, e);
        /* scaled only: the input differs from the unit mesh by one rounding per coordinate;
         * beyond the range the solver is refused */
        tg_mesh* m = transformed(sc->unit, s, 0.0);
        char how[64];
        snprintf(how, sizeof how, "x1e%d", e);
        if (s * sc->extent > 1e150) {
            CHECK_STATUS(compute(sc, m, &a), TG_ERR_UNSUPPORTED);
            tg_mesh_destroy(m);
            continue;
        }
        CHECK_STATUS(compute(sc, m, &a), TG_OK);
        compare(sc, &a, nv, s, 0.0, e, how);
        tg_mesh_destroy(m);
        sc->variants++;
        /* and moved 2^10 sizes away (its largest coordinate s * 4 * 2^10 * size must stay within
         * the range): coordinates up to 2^12 sizes are rounded by up to 2^-41 sizes, which moves
         * a distance by a few times that: allowed 2^-38 sizes beyond the relative 1e-12 */
        double t = ldexp(sc->size, 10);
        if (s * 4.0 * (t + sc->size) > 1e150) continue;
        m = transformed(sc->unit, s, t);
        snprintf(how, sizeof how, "x1e%d moved", e);
        CHECK_STATUS(compute(sc, m, &a), TG_OK);
        compare(sc, &a, nv, s, ldexp(sc->size, -38), e, how);
        tg_mesh_destroy(m);
        sc->variants++;
    }
    /* powers of two: the moved mesh scaled exactly, to the edge of the range (the unit mesh
     * moved is the reference: the same numbers up to the exponent) */
    for (int k = -490; k <= 490; k += TG_TEST_DEPTH(TG_TEST_WORK(70, 245), TG_TEST_WORK(245, 490))) {
        double s = ldexp(1.0, k);
        tg_mesh* m = transformed(sc->unit, s, ldexp(sc->size, 10));
        if (s * 4.0 * ldexp(sc->size, 11) > 1e150) {
            tg_geodesic* g = (tg_geodesic*)1;
            CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_ERR_UNSUPPORTED);
            CHECK(g == NULL);
        } else {
            char how[64];
            snprintf(how, sizeof how, "x2^%d moved", k);
            CHECK_STATUS(compute(sc, m, &a), TG_OK);
            compare(sc, &a, nv, s, 0.0, k, how); /* exact inputs */
            sc->variants++;
        }
        tg_mesh_destroy(m);
    }
    printf("%s: %d scaled or moved copies, largest relative difference %.3g (at exponent %d); %d locally shortest "
           "paths ended in another geodesic\n", sc->name, sc->variants, sc->worst, sc->worst_e, sc->other_geodesic);
    free(a.field_v), free(a.field_f), free(sc->ref.field_v), free(sc->ref.field_f);
}

/* ---- the other commands' computations at any scale ---- */

/* Everything but the field and the paths above, about spot (oded_spot_low_resolution) and the
 * same mesh scaled: farthest-point sampling (samples, distances, labels), Voronoi cells (labels,
 * distances, boundary points), isolines (points, faces, positions), a route through waypoints
 * and the distance matrix. On the mesh scaled by 2^k (k = +-330, +-490) they are the unscaled
 * results, lengths and positions times 2^k, bit for bit; at 1e100 and 1e-100 the same indices
 * and the same numbers within 1e-12 relative (positions: 1e-9 or 1e-7 of the diagonal, below).
 * These computations were scale-free before 0.5: this test guards them (it passes on the
 * code of 0.4 too) and is the table's entry for sample, field --labels,
 * field --isolines, path --through and field --sources. */
typedef struct more {
    uint32_t samples[12], *fps_label, *vor_label;
    double *fps_dist, *vor_dist, *matrix, through;
    double *curve, curve_path; /* a curve field (2 segments) and the exact path from it */
    size_t bpoints, ipoints, ipolylines;
    double *bxyz, *ixyz;
    tg_surface_point *ipts;
    uint32_t* ifaces;
} more;

static void more_compute(const tg_mesh* m, double s, more* r)
{
    size_t n = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    r->fps_label = malloc(n * sizeof *r->fps_label), r->vor_label = malloc(n * sizeof *r->vor_label);
    r->fps_dist = malloc(n * sizeof *r->fps_dist), r->vor_dist = malloc(n * sizeof *r->vor_dist);
    r->matrix = malloc(3 * n * sizeof *r->matrix);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, 12, NULL, r->samples, r->fps_dist, r->fps_label,
                                                     NULL), TG_OK);
    const tg_surface_point src[4] = {tg_surface_vertex(0), tg_surface_vertex(300), tg_surface_face(77, 0.2, 0.3, 0.5),
                                     tg_surface_edge(301, 0.37)};
    tg_voronoi_boundaries* b = NULL;
    CHECK_STATUS(tg_voronoi_boundaries_create(NULL, &b), TG_OK);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, src, 4, NULL, b, r->vor_dist, r->vor_label, NULL), TG_OK);
    tg_voronoi_boundaries_view bv;
    tg_voronoi_boundaries_get_view(b, &bv);
    r->bpoints = bv.point_count;
    r->bxyz = malloc(3 * (bv.point_count + 1) * sizeof *r->bxyz);
    memcpy(r->bxyz, bv.xyz, 3 * bv.point_count * sizeof *r->bxyz);
    tg_voronoi_boundaries_destroy(b);
    const double levels[3] = {0.1 * s, 0.35 * s, 0.6 * s};
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(g, NULL, src, 1, levels, 3, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_view iv;
    tg_isolines_get_view(iso, &iv);
    r->ipoints = iv.point_count, r->ipolylines = iv.polyline_count;
    r->ixyz = malloc(3 * (iv.point_count + 1) * sizeof *r->ixyz);
    r->ipts = malloc((iv.point_count + 1) * sizeof *r->ipts);
    r->ifaces = malloc((iv.point_count + 1) * sizeof *r->ifaces);
    if (iv.point_count) {
        memcpy(r->ixyz, iv.xyz, 3 * iv.point_count * sizeof *r->ixyz);
        memcpy(r->ipts, iv.points, iv.point_count * sizeof *r->ipts);
        memcpy(r->ifaces, iv.faces, iv.point_count * sizeof *r->ifaces);
    }
    tg_isolines_destroy(iso);
    tg_path* p = NULL;
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    CHECK_STATUS(tg_geodesic_path_through(g, NULL, src, 3, TG_PATH_OPEN, NULL, p, NULL), TG_OK);
    tg_path_view pv;
    tg_path_get_view(p, &pv);
    r->through = pv.length;
    tg_path_destroy(p);
    CHECK_STATUS(tg_geodesic_distance_matrix(g, src, 3, NULL, 1, r->matrix, NULL), TG_OK);
    /* curves: an edge of face 77 and a chord of face 100 */
    const uint32_t* t = tg_mesh_triangles(m);
    const tg_surface_segment seg[2] = {{tg_surface_vertex(t[3 * 77]), tg_surface_vertex(t[3 * 77 + 1])},
                                       {tg_surface_face(100, 0.6, 0.2, 0.2), tg_surface_edge(301, 0.37)}};
    r->curve = malloc(n * sizeof *r->curve);
    CHECK_STATUS(tg_geodesic_curve_field(g, NULL, NULL, 0, seg, 2, NULL, 0, NULL, NULL, r->curve, NULL), TG_OK);
    tg_surface_point to = tg_surface_vertex(200);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    CHECK_STATUS(tg_geodesic_curve_path(g, NULL, NULL, 0, seg, 2, &to, NULL, p), TG_OK);
    tg_path_get_view(p, &pv);
    r->curve_path = pv.length;
    tg_path_destroy(p);
    tg_geodesic_destroy(g);
}

static void more_free(more* r)
{
    free(r->fps_label), free(r->vor_label), free(r->fps_dist), free(r->vor_dist), free(r->matrix), free(r->curve);
    free(r->bxyz), free(r->ixyz), free(r->ipts), free(r->ifaces);
}

/* got / s against want: bit for bit when exact, else within rel (of `unit` for positions). */
static int more_off(const double* got, const double* want, size_t n, double s, bool exact, double rel, double unit)
{
    int off = 0;
    for (size_t i = 0; i < n; ++i) {
        if (exact) off += !(got[i] == want[i] * s) && !(isinf(got[i]) && got[i] == want[i]);
        else off += !(fabs(got[i] / s - want[i]) <= rel * (unit > 0.0 ? unit : fabs(want[i]))) && !(isinf(got[i]) && got[i] == want[i]);
    }
    return off;
}

static void test_more_commands(void)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/oded_spot_low_resolution.obj", tg_test_meshes_dir());
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &m), TG_OK);
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double diag = 0.0;
    for (int k = 0; k < 3; ++k) diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    diag = sqrt(diag);
    more ref;
    more_compute(m, 1.0, &ref);
    const double scales[] = {ldexp(1.0, -490), ldexp(1.0, -330), ldexp(1.0, 330), ldexp(1.0, 490), 1e100, 1e-100};
    for (int i = 0; i < 6; ++i) {
        double s = scales[i];
        bool exact = i < 4;
        tg_mesh* ms = transformed(m, s, 0.0);
        more r;
        more_compute(ms, s, &r);
        int idx = memcmp(r.samples, ref.samples, sizeof r.samples) != 0;
        idx += memcmp(r.fps_label, ref.fps_label, n * sizeof *r.fps_label) != 0;
        idx += memcmp(r.vor_label, ref.vor_label, n * sizeof *r.vor_label) != 0;
        idx += r.bpoints != ref.bpoints || r.ipoints != ref.ipoints || r.ipolylines != ref.ipolylines;
        if (exact && !idx && r.ipoints)
            idx += memcmp(r.ipts, ref.ipts, r.ipoints * sizeof *r.ipts) != 0 || memcmp(r.ifaces, ref.ifaces, r.ipoints * sizeof *r.ifaces) != 0;
        int num = more_off(r.fps_dist, ref.fps_dist, n, s, exact, 1e-12, 0.0) + more_off(r.vor_dist, ref.vor_dist, n, s, exact, 1e-12, 0.0) +
                  more_off(r.matrix, ref.matrix, 3 * n, s, exact, 1e-12, 0.0) + more_off(&r.through, &ref.through, 1, s, exact, 1e-12, 0.0) +
                  more_off(r.curve, ref.curve, n, s, exact, 1e-12, 0.0) + more_off(&r.curve_path, &ref.curve_path, 1, s, exact, 1e-12, 0.0);
        /* boundary crossings are found to 1e-10 (tg_geodesic_voronoi): held to 1e-9; isoline points
         * move by up to 3.3e-8 of the diagonal when the mesh is scaled by 1 + 2^-50 or by 3 (a
         * rounding of the input: points where two circles meet nearly tangentially are known to
         * about the square root of the rounding), as at 1e+-100: held to 1e-7 there */
        if (!idx)
            num += more_off(r.bxyz, ref.bxyz, 3 * r.bpoints, s, exact, 1e-9, diag) +
                   more_off(r.ixyz, ref.ixyz, 3 * r.ipoints, s, exact, 1e-7, diag);
        printf("other commands at x%g: %d index arrays and %d numbers differ (%zu samples/labels, %zu boundary and %zu "
               "isoline points, a route, a 3-row matrix, a curve field and path)\n", s, idx, num, 12 + 2 * n, r.bpoints,
               r.ipoints);
        CHECK_MSG(idx == 0 && num == 0, "x%g: %d index arrays and %d numbers differ from the unscaled ones", s, idx, num);
        more_free(&r);
        tg_mesh_destroy(ms);
    }
    more_free(&ref);
    tg_mesh_destroy(m);
}

int main(void)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/nvd_spot.obj", tg_test_meshes_dir());
    tg_mesh* spot = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &spot), TG_OK);
    tg_mesh* holed = make_plate(12, 3, 1.0);
    if (!spot || !holed) return tg_test_finish();
    static scene scenes[2];
    scenes[0].name = "spot", scenes[1].name = "holed plate";
    scenes[1].tied = true;
    scenes[0].unit = quantized(spot, &scenes[0].size, &scenes[0].extent);
    scenes[1].unit = quantized(holed, &scenes[1].size, &scenes[1].extent);
    for (int i = 0; i < 2; ++i) {
        pick_points(&scenes[i], 20261125u + (uint64_t)i);
        run_scene(&scenes[i]);
        tg_mesh_destroy(scenes[i].unit);
    }
    tg_mesh_destroy(spot);
    tg_mesh_destroy(holed);
    test_more_commands();
    return tg_test_finish();
}
