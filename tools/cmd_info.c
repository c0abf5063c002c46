/* cmd_info.c - `trigeo info MESH [--json]`: the mesh validation report. */
#include "cli.h"

#include <string.h>

static void print_json(const char* path, const tg_mesh_report* r)
{
    printf("{\n  \"file\": \"");
    for (const char* p = path; *p; ++p) {
        if (*p == '"' || *p == '\\') putchar('\\');
        if ((unsigned char)*p < 0x20) printf("\\u%04x", (unsigned char)*p);
        else putchar(*p);
    }
    printf("\",\n");
    printf("  \"vertices\": %llu,\n", (unsigned long long)r->vertices);
    printf("  \"faces\": %llu,\n", (unsigned long long)r->faces);
    printf("  \"edges\": %llu,\n", (unsigned long long)r->edges);
    printf("  \"components\": %llu,\n", (unsigned long long)r->components);
    printf("  \"boundary_edges\": %llu,\n", (unsigned long long)r->boundary_edges);
    printf("  \"boundary_loops\": %llu,\n", (unsigned long long)r->boundary_loops);
    printf("  \"nonmanifold_edges\": %llu,\n", (unsigned long long)r->nonmanifold_edges);
    printf("  \"nonmanifold_vertices\": %llu,\n", (unsigned long long)r->nonmanifold_vertices);
    printf("  \"misoriented_edges\": %llu,\n", (unsigned long long)r->misoriented_edges);
    printf("  \"degenerate_faces\": %llu,\n", (unsigned long long)r->degenerate_faces);
    printf("  \"duplicate_faces\": %llu,\n", (unsigned long long)r->duplicate_faces);
    printf("  \"unreferenced_vertices\": %llu,\n", (unsigned long long)r->unreferenced_vertices);
    printf("  \"euler_characteristic\": %lld,\n", (long long)r->euler_characteristic);
    printf("  \"closed_manifold\": %s,\n", r->closed_manifold ? "true" : "false");
    if (r->genus >= 0)
        printf("  \"genus\": %lld,\n", (long long)r->genus);
    else
        printf("  \"genus\": null,\n");
    printf("  \"bbox_min\": [%.17g, %.17g, %.17g],\n", r->bbox_min[0], r->bbox_min[1], r->bbox_min[2]);
    printf("  \"bbox_max\": [%.17g, %.17g, %.17g]\n}\n", r->bbox_max[0], r->bbox_max[1], r->bbox_max[2]);
}

static void print_text(const char* path, const tg_mesh_report* r, size_t bytes)
{
    printf("%s\n", path);
    printf("  vertices               %llu\n", (unsigned long long)r->vertices);
    printf("  faces                  %llu\n", (unsigned long long)r->faces);
    printf("  edges                  %llu\n", (unsigned long long)r->edges);
    printf("  components             %llu\n", (unsigned long long)r->components);
    printf("  boundary edges         %llu in %llu loop(s)\n", (unsigned long long)r->boundary_edges,
           (unsigned long long)r->boundary_loops);
    printf("  non-manifold edges     %llu\n", (unsigned long long)r->nonmanifold_edges);
    printf("  non-manifold vertices  %llu\n", (unsigned long long)r->nonmanifold_vertices);
    printf("  misoriented edges      %llu\n", (unsigned long long)r->misoriented_edges);
    printf("  degenerate faces       %llu\n", (unsigned long long)r->degenerate_faces);
    printf("  duplicate faces        %llu\n", (unsigned long long)r->duplicate_faces);
    printf("  unreferenced vertices  %llu\n", (unsigned long long)r->unreferenced_vertices);
    printf("  Euler characteristic   %lld\n", (long long)r->euler_characteristic);
    if (r->genus >= 0)
        printf("  genus                  %lld (closed manifold)\n", (long long)r->genus);
    else
        printf("  genus                  n/a (%s)\n", r->closed_manifold ? "non-orientable" : "not a closed manifold");
    printf("  bounding box           [%.6g, %.6g, %.6g] - [%.6g, %.6g, %.6g]\n", r->bbox_min[0],
           r->bbox_min[1], r->bbox_min[2], r->bbox_max[0], r->bbox_max[1], r->bbox_max[2]);
    printf("  memory                 %.1f MiB (%.1f bytes/face)\n", bytes / 1048576.0,
           r->faces ? (double)bytes / (double)r->faces : 0.0);
}

static int run(int argc, char** argv)
{
    const char* path = NULL;
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--json"))
            json = true;
        else if (argv[i][0] == '-' && argv[i][1])
            return cli_usage("info", "unknown option '%s'", argv[i]);
        else if (!path)
            path = argv[i];
        else
            return cli_usage("info", "unexpected argument '%s'", argv[i]);
    }
    if (!path) return cli_usage("info", "missing MESH");
    tg_mesh* mesh = cli_load_mesh(path);
    if (!mesh) return CLI_INPUT;
    const tg_mesh_report* r = tg_mesh_get_report(mesh);
    if (json)
        print_json(path, r);
    else
        print_text(path, r, tg_mesh_memory_bytes(mesh));
    tg_mesh_destroy(mesh);
    return CLI_OK;
}

const cli_command cli_cmd_info = {
    "info", "info MESH [--json]",
    "Loads MESH and prints its validation report: counts of vertices, faces, edges, components,\n"
    "boundary edges and loops, non-manifold edges and (pinched) vertices, inconsistently oriented\n"
    "edges, degenerate (zero-area) and duplicate faces, unreferenced vertices, the Euler\n"
    "characteristic, the genus when the mesh is a closed manifold, and the bounding box.\n\n"
    "  --json   machine-readable output; genus is null when not a closed manifold\n",
    run,
};
