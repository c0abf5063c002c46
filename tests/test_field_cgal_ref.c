/* test_field_cgal_ref.c - exact fields against an independent exact implementation: CGAL's
 * Surface_mesh_shortest_path (Xin & Wang's window propagation, exact predicates), whose distances
 * for a vertex, a face point 1e-3 from an edge and a face point source on 11 corpus meshes (scans,
 * CAD, open surfaces with holes, genus 3) are committed in tests/ref/ with the script that made
 * them (tests/ref/make_field_refs.sh). Sources exactly on an edge are not compared: CGAL 5.5
 * misplaces them (its distance to an end vertex of the source's own edge comes out below the
 * Euclidean distance); they are checked by symmetry (test_field_engine) and known answers. Every reference vertex must agree within 1e-12 of the field's
 * largest distance, inf where CGAL finds no path. The exact paths from each source to 20 of the
 * reference vertices must have CGAL's length within 1e-9 relative, be proven and certified.
 * The default method (options all zero, and NULL options) on the same fixed pairs: the share of
 * globally shortest paths (CGAL's length within 1e-9 relative) must be at least 98%, and every
 * path it labels proven must be globally shortest. The other methods on the
 * first pairs: valid paths (tg_test_path.h), never shorter than CGAL's distance. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"
#include "tg_test_path.h"

typedef tg_test_ref_entry entry;

/* The default method's record over every pair of every file: [0] all-zero options, [1] NULL. */
typedef struct default_tally {
    size_t pairs, shortest, proven;
} default_tally;
static default_tally default_tallies[2];

/* The default method is globally shortest on at least this share of random pairs. */
#define DEFAULT_SHORTEST_SHARE 0.98

/* One pair through the default method, both ways of asking for it: tallied, and a path labelled
 * proven must have CGAL's length within 1e-9 relative (the label's promise). */
static void tally_default(const char* file, const char* spec, tg_geodesic* g, tg_geodesic_workspace* ws,
                          const tg_surface_point* s, const entry* e, tg_path* path)
{
    tg_path_options zero;
    memset(&zero, 0, sizeof zero);
    tg_surface_point t = tg_surface_vertex(e->v);
    for (int k = 0; k < 2; ++k) {
        CHECK_STATUS(tg_geodesic_path(g, ws, s, &t, k ? NULL : &zero, path), TG_OK);
        tg_path_view v;
        tg_path_get_view(path, &v);
        bool shortest = fabs(v.length - e->d) <= 1e-9 * e->d;
        default_tally* d = &default_tallies[k];
        d->pairs++;
        d->shortest += shortest;
        if (v.global != TG_PATH_PROVEN) continue;
        d->proven++;
        CHECK_MSG(shortest, "%s %s -> v:%u: the default (%s options) labelled proven a path of %.17g, CGAL %.17g", file,
                  spec, e->v, k ? "NULL" : "zero", v.length, e->d);
    }
}

/* Exact paths (TG_PATH_EXACT) from the source to the first reference vertices: the length is
 * CGAL's distance within 1e-9 relative (never shorter beyond rounding), the path is proven and
 * certified straight: an independent exact reference for paths. */
static void compare_paths(const char* file, const tg_mesh* m, tg_geodesic* g, const char* spec,
                          const tg_surface_point* s, const entry* e, size_t n, double far)
{
    tg_geodesic_workspace* ws = NULL;
    tg_path* path = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &path), TG_OK);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = TG_PATH_EXACT;
    /* exact paths a source: 20 in the full suite (4 under the sanitizers), 6 (3) in the fast one */
    size_t count = 0, want = TG_TEST_DEPTH(TG_TEST_WORK(20, 4), TG_TEST_WORK(6, 3));
    double worst = 0.0, cert = 0.0;
    for (size_t i = 0; i < n && count < want && ws && path; ++i) {
        if (!isfinite(e[i].d) || e[i].d < 1e-6 * far) continue; /* unreachable, or at the source */
        tg_surface_point t = tg_surface_vertex(e[i].v);
        CHECK_STATUS(tg_geodesic_path(g, ws, s, &t, &o, path), TG_OK);
        tg_path_view v;
        tg_path_get_view(path, &v);
        double rel = (v.length - e[i].d) / e[i].d;
        if (fabs(rel) > worst) worst = fabs(rel);
        if (v.max_angle_defect > cert) cert = v.max_angle_defect;
        CHECK_MSG(fabs(rel) <= 1e-9 && v.global == TG_PATH_PROVEN && v.max_angle_defect <= 1e-10,
                  "%s %s -> v:%u: exact path %.17g (%s, certificate %.2g), CGAL %.17g", file, spec, e[i].v, v.length,
                  tg_path_global_name(v.global), v.max_angle_defect, e[i].d);
        tally_default(file, spec, g, ws, s, &e[i], path);
        /* the local methods: valid paths, never shorter than the distance (the slow relaxation on
         * one pair of the smaller meshes) */
        for (int k = 1; k < 4 && count < TG_TEST_WORK(5, 2); ++k) {
            tg_path_options lo;
            memset(&lo, 0, sizeof lo);
            lo.method = tg_test_path_methods[k];
            if (lo.method == TG_PATH_RELAX && (count > 0 || tg_mesh_face_count(m) > 8000)) continue;
            CHECK_STATUS(tg_geodesic_path(g, ws, s, &t, &lo, path), TG_OK);
            tg_path_get_view(path, &v);
            tg_test_check_path(tg_test_method_name(lo.method), m, &v, s, &t, 0);
            CHECK_MSG(v.length >= e[i].d * (1 - 1e-9), "%s %s -> v:%u: %s path %.17g below CGAL's %.17g", file, spec,
                      e[i].v, tg_test_method_name(lo.method), v.length, e[i].d);
        }
        count++;
    }
    CHECK_MSG(count == want, "%s %s: only %zu reachable reference vertices for paths", file, spec, count);
    printf("%s %s: %zu exact paths, largest relative difference %.2g, largest certificate %.2g rad\n", file, spec, count,
           worst, cert);
    tg_path_destroy(path);
    tg_geodesic_workspace_destroy(ws);
}

/* Compares the field of one source with its reference entries. */
static void compare(const char* file, const tg_mesh* m, tg_geodesic* g, const char* spec, const entry* e, size_t n)
{
    size_t nv = tg_mesh_vertex_count(m);
    tg_surface_point s;
    if (!tg_test_parse_spec(spec, &s)) {
        CHECK_MSG(0, "%s: bad source '%s'", file, spec);
        return;
    }
    double* d = malloc(nv * sizeof *d);
    CHECK_STATUS(tg_geodesic_field(g, NULL, &s, 1, NULL, d, NULL), TG_OK);
    double far = 0, worst = 0;
    for (size_t i = 0; i < n; ++i)
        if (isfinite(e[i].d) && e[i].d > far) far = e[i].d;
    size_t at = 0;
    for (size_t i = 0; i < n; ++i) {
        CHECK(e[i].v < nv);
        if (e[i].v >= nv) break;
        double ours = d[e[i].v];
        if (isinf(e[i].d) || isinf(ours)) {
            CHECK_MSG(isinf(e[i].d) && isinf(ours), "%s %s: vertex %u: trigeo %.17g, CGAL %.17g", file, spec, e[i].v, ours,
                      e[i].d);
            continue;
        }
        double diff = fabs(ours - e[i].d);
        if (diff > worst) worst = diff, at = i;
    }
    CHECK_MSG(worst <= 1e-12 * far, "%s %s: vertex %u: trigeo %.17g, CGAL %.17g (%.2g of the largest distance)", file, spec,
              e[at].v, d[e[at].v], e[at].d, far > 0 ? worst / far : 0.0);
    printf("%s %s: %zu vertices, largest difference %.2g of the largest distance %.6g\n", file, spec, n,
           far > 0 ? worst / far : 0.0, far);
    free(d);
    compare_paths(file, m, g, spec, &s, e, n, far);
}

/* The mesh of the reference file being read and its solver, made when its "mesh" line is seen. */
typedef struct ref_state {
    char mesh[256];
    tg_mesh* m;
    tg_geodesic* g;
} ref_state;

static void each_source(const char* mesh_file, const char* spec, const tg_test_ref_entry* e, size_t n, void* ctx)
{
    ref_state* st = (ref_state*)ctx;
    if (strcmp(st->mesh, mesh_file) != 0) {
        tg_geodesic_destroy(st->g), tg_mesh_destroy(st->m);
        st->g = NULL;
        snprintf(st->mesh, sizeof st->mesh, "%s", mesh_file);
        st->m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), mesh_file);
        if (st->m) CHECK_STATUS(tg_geodesic_create(st->m, NULL, &st->g), TG_OK);
    }
    if (st->g) compare(mesh_file, st->m, st->g, spec, e, n);
}

static void check_file(const char* name)
{
    ref_state st;
    memset(&st, 0, sizeof st);
    int sources = tg_test_read_ref(name, each_source, &st);
    CHECK_MSG(sources == 3, "%s: %d sources", name, sources);
    tg_geodesic_destroy(st.g);
    tg_mesh_destroy(st.m);
}

int main(void)
{
    const char* files[] = {"nvd_spot", "igl_bunny", "cgal_fandisk", "cgal_elephant-with-holes", "oded_plane_holes",
                           "igl_decimated-knight", "cgal_pinion", "igl_3holes", "lpm_blub_triangulated", "cgal_turbine",
                           "c3d_teapot"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) check_file(files[i]);
    for (int k = 0; k < 2; ++k) {
        const default_tally* d = &default_tallies[k];
        double share = d->pairs ? (double)d->shortest / (double)d->pairs : 0.0;
        printf("default method (%s options): %zu of %zu pairs globally shortest (%.2f%%), %zu labelled proven\n",
               k ? "NULL" : "zero", d->shortest, d->pairs, 100.0 * share, d->proven);
        CHECK_MSG(d->pairs > 0 && share >= DEFAULT_SHORTEST_SHARE,
                  "default method (%s options): globally shortest on %.2f%% of %zu pairs, below %.0f%%", k ? "NULL" : "zero",
                  100.0 * share, d->pairs, 100.0 * DEFAULT_SHORTEST_SHARE);
    }
    return tg_test_finish();
}
