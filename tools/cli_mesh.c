/* cli_mesh.c - the mesh of a command: read from a file or standard input in the format that
 * --format names (else the file's extension or content), the reader's warnings printed, and for
 * distances coordinates beyond the range where squared distances stay finite refused.
 * Based on: the CLI contract of the project's DESIGN.md (inputs, error format). */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* --format of the command line (any command): the mesh's format instead of its extension. */
static tg_format mesh_format = TG_FORMAT_AUTO;

void cli_set_mesh_format(tg_format format) { mesh_format = format; }

tg_mesh* cli_load_mesh(const char* path)
{
    tg_diag diag;
    tg_mesh* mesh = NULL;
    tg_status st;
    if (!strcmp(path, "-")) {
        size_t n = 0;
        char* data = cli_read_all("-", &n);
        if (!data) return NULL;
        st = tg_mesh_load_memory(data, n, "-", mesh_format, NULL, &diag, &mesh);
        free(data);
    } else {
        st = tg_mesh_load(path, mesh_format, NULL, &diag, &mesh);
    }
    if (st != TG_OK) {
        cli_error_diag(&diag, st);
        return NULL;
    }
    if (diag.message[0]) cli_error_diag(&diag, st); /* a warning: something the reader tolerated */
    return mesh;
}

tg_mesh* cli_load_mesh_for_distances(const char* path)
{
    tg_mesh* m = cli_load_mesh(path);
    if (!m) return NULL;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    for (int k = 0; k < 3; ++k)
        if (tg_mesh_vertex_count(m) && !(r->bbox_min[k] >= -1e150 && r->bbox_max[k] <= 1e150)) {
            cli_error(path, 0,
                      "coordinates reach %s, beyond the supported range of +-1e150 for distances (squared "
                      "distances would overflow): rescale the mesh",
                      cli_num(fabs(r->bbox_min[k]) > fabs(r->bbox_max[k]) ? r->bbox_min[k] : r->bbox_max[k]).s);
            tg_mesh_destroy(m);
            return NULL;
        }
    return m;
}
