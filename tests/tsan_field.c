/* tsan_field.c - the driver of cli_tsan_field.sh: one field on 2, 3 and 7 threads (the crew and
 * its lanes), built with the library's sources under ThreadSanitizer; exit 1 when two thread
 * counts disagree. usage: tsan_field MESH... */
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
        printf("%s: %zu vertices on 2, 3 and 7 threads\n", argv[a], n);
        free(ref), free(got);
        tg_geodesic_destroy(g);
        tg_mesh_destroy(m);
    }
    return bad;
}
