/* tsan_field.c - the driver of cli_tsan_field.sh: one field on 2, 3 and 7 threads (the crew and
 * its lanes), and the calls whose lanes carry more (points, the log map's records, isolines'
 * recorded windows) on 2 and 7, built with the library's sources under ThreadSanitizer; exit 1
 * when two thread counts disagree. usage: tsan_field MESH... */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

int main(int argc, char** argv)
{
    int bad = 0;
    for (int a = 1; a < argc; ++a) {
        tg_mesh* m = NULL;
        tg_diag d;
        tg_geodesic* g = NULL;
        if (tg_mesh_load(argv[a], TG_FORMAT_AUTO, NULL, &d, &m) != TG_OK || tg_geodesic_create(m, NULL, &g) != TG_OK) {
            fprintf(stderr, "tsan_field: cannot load %s\n", argv[a]);
            return 2;
        }
        size_t n = tg_mesh_vertex_count(m);
        double *ref = malloc(n * sizeof *ref), *got = malloc(n * sizeof *got);
        tg_surface_point s[2] = {tg_surface_vertex(0), tg_surface_face(0, 0.2, 0.3, 0.5)};
        static const int counts[3] = {2, 3, 7};
        for (int k = 0; k < 3; ++k) {
            tg_field_options o;
            memset(&o, 0, sizeof o);
            o.threads = counts[k];
            if (tg_geodesic_field(g, NULL, s, 2, &o, k ? got : ref, NULL) != TG_OK) bad = 1;
            if (k && memcmp(ref, got, n * sizeof *ref)) {
                fprintf(stderr, "tsan_field: %s: %d threads differ from 2\n", argv[a], counts[k]);
                bad = 1;
            }
        }
        /* points, log map, isolines: 2 and 7 threads */
        double *ang[2], at[2][4], lv = 0.5 * ref[n / 2];
        tg_surface_point pts[4] = {tg_surface_vertex((uint32_t)(n / 2)), tg_surface_face(1, 0.3, 0.3, 0.4),
                                   tg_surface_face((uint32_t)(tg_mesh_face_count(m) / 2), 0.1, 0.1, 0.8),
                                   tg_surface_edge(3, 0.5)};
        size_t iso_points[2] = {0, 0};
        for (int k = 0; k < 2; ++k) {
            tg_field_options o;
            memset(&o, 0, sizeof o);
            o.threads = k ? 7 : 2;
            ang[k] = malloc(n * sizeof(double));
            if (tg_geodesic_log_map(g, NULL, s + 1, NULL, &o, k ? got : ref, ang[k], NULL) != TG_OK) bad = 1;
            if (tg_geodesic_field_at(g, NULL, s, 1, pts, 4, &o, at[k], NULL, NULL) != TG_OK) bad = 1;
            tg_isolines* iso = NULL;
            tg_isolines_view v;
            if (tg_isolines_create(NULL, &iso) != TG_OK || !(lv > 0.0) ||
                tg_geodesic_isolines(g, NULL, s, 1, &lv, 1, &o, iso, NULL, NULL) != TG_OK)
                bad = 1;
            tg_isolines_get_view(iso, &v);
            iso_points[k] = v.point_count;
            tg_isolines_destroy(iso);
        }
        if (memcmp(ref, got, n * sizeof *ref) || memcmp(ang[0], ang[1], n * sizeof(double)) ||
            memcmp(at[0], at[1], sizeof at[0]) || iso_points[0] != iso_points[1] || !iso_points[0]) {
            fprintf(stderr, "tsan_field: %s: the log map, points or isolines differ on 2 and 7 threads\n", argv[a]);
            bad = 1;
        }
        free(ang[0]), free(ang[1]);
        printf("%s: %zu vertices on 2, 3 and 7 threads; log map, points, isolines (%zu points) on 2 and 7\n",
               argv[a], n, iso_points[0]);
        free(ref), free(got);
        tg_geodesic_destroy(g);
        tg_mesh_destroy(m);
    }
    return bad;
}
